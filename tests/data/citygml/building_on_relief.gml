<?xml version="1.0" encoding="UTF-8"?>
<!-- CityGML 2.0 for tests/geometry/CityGmlTest.cpp: a LoD1 building on a TIN relief of two
     triangles (sloping from 10 m at x = 0 to 20 m at x = 100), and a tree (an ignored type). -->
<CityModel xmlns="http://www.opengis.net/citygml/2.0" xmlns:bldg="http://www.opengis.net/citygml/building/2.0" xmlns:dem="http://www.opengis.net/citygml/relief/2.0" xmlns:veg="http://www.opengis.net/citygml/vegetation/2.0" xmlns:gml="http://www.opengis.net/gml">
  <gml:boundedBy><gml:Envelope srsName="EPSG:28992" srsDimension="3"/></gml:boundedBy>
  <cityObjectMember>
    <dem:ReliefFeature gml:id="relief">
      <dem:lod>1</dem:lod>
      <dem:reliefComponent>
        <dem:TINRelief gml:id="tin">
          <dem:lod>1</dem:lod>
          <dem:tin><gml:TriangulatedSurface><gml:trianglePatches>
            <gml:Triangle><gml:exterior><gml:LinearRing><gml:posList>0 0 10 100 0 20 100 100 20 0 0 10</gml:posList></gml:LinearRing></gml:exterior></gml:Triangle>
            <gml:Triangle><gml:exterior><gml:LinearRing><gml:posList>0 0 10 100 100 20 0 100 10 0 0 10</gml:posList></gml:LinearRing></gml:exterior></gml:Triangle>
          </gml:trianglePatches></gml:TriangulatedSurface></dem:tin>
        </dem:TINRelief>
      </dem:reliefComponent>
    </dem:ReliefFeature>
  </cityObjectMember>
  <cityObjectMember>
    <veg:SolitaryVegetationObject gml:id="tree">
      <veg:lod1Geometry><gml:MultiSurface><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing>
        <gml:posList>70 70 15 72 70 15 72 72 15 70 70 15</gml:posList>
      </gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></veg:lod1Geometry>
    </veg:SolitaryVegetationObject>
  </cityObjectMember>
  <cityObjectMember>
    <bldg:Building gml:id="house">
      <bldg:lod1MultiSurface><gml:MultiSurface>
        <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>40 40 14 40 50 14 50 50 14 50 40 14 40 40 14</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
        <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>40 40 24 50 40 24 50 50 24 40 50 24 40 40 24</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
        <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>40 40 14 50 40 14 50 40 24 40 40 24 40 40 14</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
        <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>50 40 14 50 50 14 50 50 24 50 40 24 50 40 14</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
        <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>50 50 14 40 50 14 40 50 24 50 50 24 50 50 14</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
        <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>40 50 14 40 40 14 40 40 24 40 50 24 40 50 14</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
      </gml:MultiSurface></bldg:lod1MultiSurface>
    </bldg:Building>
  </cityObjectMember>
</CityModel>
